//! u-blox UBX frames: the framing layer (spec/binary/ubx/protocol.yaml) and what the generated
//! messages (`nmeaspec::ubx_messages`) read and write their payloads with.
//!
//! The Rust side of the Python runtime's ubx.py, with its rules and error messages. A frame is the
//! sync bytes B5 62, a class and an id byte, the payload's length (two bytes, little endian) and
//! the payload, closed by a Fletcher-8 checksum over class to payload. Decoding reads the payload
//! in place and allocates nothing: characters, bytes, a repeated group's entries and the bytes
//! after a layout are views of the payload. Encoding writes the whole frame into a caller's
//! buffer. What a decoder keeps as sent (reserved bytes, the bits of a bitfield no part names, a
//! NaN's bits, bytes after the layout) is written back as it was. Facts from u-blox UBX-13003221
//! (u-blox 8 / M8 Receiver description, "UBX protocol": frame structure and checksum).

use core::fmt::{self, Write};
use core::marker::PhantomData;

use super::ais::JsonObject;
use super::stream::{FrameFormat, Protocol};

/// The two sync bytes every frame starts with.
pub const SYNC: [u8; 2] = [0xB5, 0x62];
/// Sync, class, id and length.
pub const HEADER_SIZE: usize = 6;
/// The two checksum bytes closing a frame.
pub const CHECKSUM_SIZE: usize = 2;
/// The most bytes a payload holds (its length field's largest value).
pub const MAX_PAYLOAD: usize = 0xFFFF;

/// The two checksum bytes (CK_A, CK_B) of `data`: 8-bit Fletcher, both sums modulo 256.
///
/// Eight bytes a step, as the C pair's `ubx_checksum` takes them: a 64-bit word is four 16-bit
/// lanes of its even bytes and four of its odd ones, each lane its own A (the sum of its bytes)
/// and B (the sum of A over the steps before), two steps at a time (the second's B takes the
/// first's bytes). The lanes are brought back modulo 256 (a mask, so that no lane carries into the
/// next) every 112 bytes, before a B could outgrow 16 bits. The bytes after the last whole step are
/// the last eight bytes' word shifted down: a step of those bytes after `pad` zeros, which add
/// nothing to A and `pad` times A to B, taken off at the end. A is then the lanes' sum and B eight
/// times their B plus each lane's A weighted by the running sums its byte is in (8 for a step's
/// first byte, ..., 1 for its last), each a weighted sum of lanes read as the top lane of a
/// product. No chain of one addition a byte: about a fifth of the byte loop's time on a frame of 50
/// bytes. Under eight bytes, byte by byte.
pub fn fletcher8(data: &[u8]) -> [u8; 2] {
    const LANES: u64 = 0x00FF_00FF_00FF_00FF;
    let word = |bytes: &[u8]| u64::from_le_bytes(bytes.try_into().unwrap_or([0; 8]));
    if data.len() < 8 {
        let (mut a, mut b) = (0u8, 0u8);
        for &byte in data {
            a = a.wrapping_add(byte);
            b = b.wrapping_add(a);
        }
        return [a, b];
    }
    // (even, odd, before) after one step of word `w`
    let step = |(even, odd, before): (u64, u64, u64), w: u64| {
        ((even + (w & LANES)) & LANES, (odd + (w >> 8 & LANES)) & LANES, (before + even + odd) & LANES)
    };
    let (mut even, mut odd, mut before) = (0u64, 0u64, 0u64);
    let mut rest = data;
    while rest.len() >= 16 {
        let (block, tail) = rest.split_at(if rest.len() >= 112 { 112 } else { rest.len() & !15 });
        let (mut e, mut o, mut b) = (even, odd, before);
        for pair in block.chunks_exact(16) {
            let (w, v) = (word(&pair[..8]), word(&pair[8..]));
            b += 2 * (e + o) + (w & LANES) + (w >> 8 & LANES);
            e += (w & LANES) + (v & LANES);
            o += (w >> 8 & LANES) + (v >> 8 & LANES);
        }
        (even, odd, before) = (e & LANES, o & LANES, b & LANES);
        rest = tail;
    }
    if rest.len() >= 8 {
        (even, odd, before) = step((even, odd, before), word(&rest[..8]));
        rest = &rest[8..];
    }
    let pad = (8 - rest.len() as u64) % 8;
    if !rest.is_empty() {
        (even, odd, before) = step((even, odd, before), word(&data[data.len() - 8..]) >> (8 * pad));
    }
    let top = |lanes: u64, weights: u64| lanes.wrapping_mul(weights) >> 48;
    let a = top(even + odd, 0x0001_0001_0001_0001);
    let b = (8 * top(before, 0x0001_0001_0001_0001))
        .wrapping_add(top(even, 0x0008_0006_0004_0002))
        .wrapping_add(top(odd, 0x0007_0005_0003_0001))
        .wrapping_sub(pad * a);
    [a as u8, b as u8]
}

/// What is wrong with a frame, a payload or a message to encode.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UbxErrorKind {
    /// The frame does not start with B5 62.
    BadSync,
    /// The frame is shorter than its header or than its length field says.
    ShortFrame,
    /// The frame is longer than its length field says.
    LongFrame,
    /// The checksum bytes are not the Fletcher-8 of class to payload.
    BadChecksum,
    /// The payload ends before a field's last byte (or a group's last entry).
    ShortPayload,
    /// A value to encode its field cannot hold (characters or bytes of another size).
    BadValue,
    /// The payload to encode is over 65,535 bytes, or the buffer cannot hold the frame.
    BufferTooSmall,
}

impl UbxErrorKind {
    /// The kind as the JSON contract names it.
    pub const fn as_str(self) -> &'static str {
        match self {
            UbxErrorKind::BadSync => "bad_sync",
            UbxErrorKind::ShortFrame => "short_frame",
            UbxErrorKind::LongFrame => "long_frame",
            UbxErrorKind::BadChecksum => "bad_checksum",
            UbxErrorKind::ShortPayload => "short_payload",
            UbxErrorKind::BadValue => "bad_value",
            UbxErrorKind::BufferTooSmall => "buffer_too_small",
        }
    }
}

/// The facts an error message is written from (`CheckEnd`: another protocol's checksum and end
/// bytes, as big-endian numbers of `width` bytes).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Detail {
    Sync { expected: [u8; 3], want: usize, sent: [u8; 3], len: usize },
    Header { need: usize, have: usize },
    Length { size: usize, have: usize },
    Checksum { sent: [u8; 2], computed: [u8; 2] },
    CheckEnd { sent: u32, computed: u32, width: usize },
    Short { offset: usize, width: usize, length: usize },
    FewEntries { count: usize, at_least: bool, width: usize, left: usize },
    Stride { stride: usize, group: &'static str, width: usize },
    StrideWritten { written: usize, group: &'static str, stride: usize },
    Size { expected: usize, found: usize },
    Buffer { need: usize, have: usize },
}

/// A UBX error (or one of another binary protocol whose messages the spec types: SkyTraq, SiRF,
/// CASIC): its kind, the message (`NAV-PVT`, or `0x01 0x07` before a layout names it) and the
/// field it concerns when known.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct UbxError {
    /// What is wrong.
    pub kind: UbxErrorKind,
    /// The protocol as errors name it: `UBX`, `SKYTRAQ`, `SIRF`, `CASIC`.
    pub protocol: &'static str,
    /// The message's name (`NAV-PVT`); empty before the frame's class and id are read.
    pub message: &'static str,
    /// The class and id of the frame, once read.
    pub class_id: Option<(u8, u8)>,
    /// The field being read or written.
    pub field: Option<&'static str>,
    detail: Detail,
}

impl UbxError {
    fn frame(kind: UbxErrorKind, class_id: Option<(u8, u8)>, detail: Detail) -> Self {
        UbxError { kind, protocol: "UBX", message: "", class_id, field: None, detail }
    }

    /// The error's address as the Python runtime gives it: `UBX NAV-PVT`, `UBX 0x01 0x07`, `UBX`.
    pub fn address(&self) -> impl fmt::Display + '_ {
        Address(self)
    }

    /// The error's message alone (`"lat needs bytes 28-31, the payload has 28"`).
    pub fn text(&self) -> impl fmt::Display + '_ {
        Message(self)
    }

    /// The error as the tools' JSON error object (the Python runtime's `error_json`): its kind,
    /// its address (`UBX NAV-PVT`), the field at fault as its name, and its message.
    pub fn write_json<W: Write + ?Sized>(&self, w: &mut W) -> fmt::Result {
        write!(w, "{{\"kind\":\"{}\",\"address\":\"{}\",\"field\":null,\"name\":", self.kind.as_str(), self.address())?;
        match self.field {
            Some(field) => write!(w, "\"{field}\"")?,
            None => w.write_str("null")?,
        }
        w.write_str(",\"message\":")?;
        super::write::write_json_display(w, &self.text())?;
        w.write_char('}')
    }
}

struct Address<'e>(&'e UbxError);

impl fmt::Display for Address<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.0.protocol)?;
        match (self.0.message, self.0.class_id) {
            ("", Some((class, id))) => write!(f, " 0x{class:02X} 0x{id:02X}"),
            ("", None) => Ok(()),
            (name, _) => write!(f, " {name}"),
        }
    }
}

struct Message<'e>(&'e UbxError);

impl fmt::Display for Message<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let field = self.0.field.unwrap_or("");
        match self.0.detail {
            Detail::Sync { expected, want, sent, len } => {
                write!(f, "a {} frame starts with", self.0.protocol)?;
                expected.iter().take(want).try_for_each(|byte| write!(f, " {byte:02X}"))?;
                f.write_str(", not")?;
                sent.iter().take(len).try_for_each(|byte| write!(f, " {byte:02X}"))
            }
            Detail::Header { need, have } => {
                write!(f, "a {} header needs {need} bytes, there are {have}", self.0.protocol)
            }
            Detail::Length { size, have } => write!(f, "the length field says {size} bytes, the frame has {have}"),
            Detail::Checksum { sent, computed } => {
                write!(f, "checksum {:02X} {:02X}, computed {:02X} {:02X}", sent[0], sent[1], computed[0], computed[1])
            }
            Detail::CheckEnd { sent, computed, width } => {
                f.write_str("checksum and end")?;
                (0..width).rev().try_for_each(|i| write!(f, " {:02X}", sent >> (8 * i) & 0xFF))?;
                f.write_str(", computed")?;
                (0..width).rev().try_for_each(|i| write!(f, " {:02X}", computed >> (8 * i) & 0xFF))
            }
            Detail::Short { offset, width, length } => {
                let (first, last) = (offset, offset + width - 1);
                if first == last {
                    write!(f, "{field} needs byte {first}, the payload has {length}")
                } else {
                    write!(f, "{field} needs bytes {first}-{last}, the payload has {length}")
                }
            }
            Detail::FewEntries { count, at_least, width, left } => write!(
                f,
                "{field} needs {}{count} entries of {} bits, {} bits left",
                if at_least { "at least " } else { "" },
                8 * width,
                8 * left
            ),
            Detail::Stride { stride, group, width } => {
                write!(f, "{field} is {stride}, an entry of {group} takes at least {width} bytes")
            }
            Detail::StrideWritten { written, group, stride } => {
                write!(f, "{field} takes the bytes of each entry of {group} ({written}), not {stride}")
            }
            Detail::Size { expected, found } => write!(f, "{field} takes {expected} bytes, not {found}"),
            Detail::Buffer { need, have } => write!(f, "the frame takes {need} bytes, the buffer has {have}"),
        }
    }
}

impl fmt::Display for UbxError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}: {}", self.kind.as_str(), self.address(), self.text())
    }
}

#[cfg(feature = "std")]
impl std::error::Error for UbxError {}

/// One whole frame, its sync bytes, length and checksum checked: its class, id and payload.
pub fn split_frame(data: &[u8]) -> Result<(u8, u8, &[u8]), UbxError> {
    let sync = data.len().min(2);
    if !matches!(data, [0xB5, 0x62, ..]) && data[..sync] != SYNC[..sync] {
        let mut sent = [0u8; 3];
        sent[..sync].copy_from_slice(&data[..sync]);
        let expected = [SYNC[0], SYNC[1], 0];
        return Err(UbxError::frame(UbxErrorKind::BadSync, None, Detail::Sync { expected, want: 2, sent, len: sync }));
    }
    if data.len() < HEADER_SIZE {
        return Err(UbxError::frame(
            UbxErrorKind::ShortFrame,
            None,
            Detail::Header { need: HEADER_SIZE, have: data.len() },
        ));
    }
    let class_id = Some((data[2], data[3]));
    let size = HEADER_SIZE + usize::from(u16::from_le_bytes([data[4], data[5]])) + CHECKSUM_SIZE;
    let detail = Detail::Length { size, have: data.len() };
    if data.len() < size {
        return Err(UbxError::frame(UbxErrorKind::ShortFrame, class_id, detail));
    }
    if data.len() > size {
        return Err(UbxError::frame(UbxErrorKind::LongFrame, class_id, detail));
    }
    let computed = fletcher8(&data[2..size - CHECKSUM_SIZE]);
    let sent = [data[size - 2], data[size - 1]];
    if sent != computed {
        return Err(UbxError::frame(UbxErrorKind::BadChecksum, class_id, Detail::Checksum { sent, computed }));
    }
    Ok((data[2], data[3], &data[HEADER_SIZE..size - CHECKSUM_SIZE]))
}

/// A payload's little-endian fields, read in order; errors name the message and the field.
#[derive(Clone, Debug)]
pub struct ByteReader<'a> {
    payload: &'a [u8],
    pos: usize,
    protocol: &'static str,
    message: &'static str,
    class_id: (u8, u8),
}

impl<'a> ByteReader<'a> {
    /// A reader at the start of `payload` of message `message` (`NAV-PVT`), class and id `class_id`.
    pub fn new(payload: &'a [u8], message: &'static str, class_id: (u8, u8)) -> Self {
        ByteReader { payload, pos: 0, protocol: "UBX", message, class_id }
    }

    /// The reader of a message of another protocol (`SKYTRAQ`, `SIRF`, `CASIC`), whose errors name it.
    pub fn of_protocol(self, protocol: &'static str) -> Self {
        ByteReader { protocol, ..self }
    }

    /// The bytes not read yet.
    pub fn remaining(&self) -> usize {
        self.payload.len() - self.pos
    }

    /// The bytes read so far.
    pub fn position(&self) -> usize {
        self.pos
    }

    fn error(&self, kind: UbxErrorKind, field: &'static str, detail: Detail) -> UbxError {
        UbxError {
            kind,
            protocol: self.protocol,
            message: self.message,
            class_id: Some(self.class_id),
            field: Some(field),
            detail,
        }
    }

    /// The next `width` bytes, for field `field`.
    pub fn bytes(&mut self, width: usize, field: &'static str) -> Result<&'a [u8], UbxError> {
        match self.payload.get(self.pos..self.pos + width) {
            Some(bytes) => {
                self.pos += width;
                Ok(bytes)
            }
            None => Err(self.error(
                UbxErrorKind::ShortPayload,
                field,
                Detail::Short { offset: self.pos, width, length: self.payload.len() },
            )),
        }
    }

    /// The next `N` bytes, for a number.
    pub fn array<const N: usize>(&mut self, field: &'static str) -> Result<[u8; N], UbxError> {
        let mut out = [0u8; N];
        out.copy_from_slice(self.bytes(N, field)?);
        Ok(out)
    }

    /// The next `N` bytes, those of a run of fields at fixed offsets (`fields`: each one's name and
    /// bytes, in order, `N` in all), after one length check for the whole run; a payload too short
    /// for the run names the first field it cuts, as reading field by field would.
    #[inline]
    pub fn run<const N: usize>(&mut self, fields: &[(&'static str, usize)]) -> Result<&'a [u8; N], UbxError> {
        match self.payload.get(self.pos..).and_then(<[u8]>::first_chunk::<N>) {
            Some(bytes) => {
                self.pos += N;
                Ok(bytes)
            }
            None => Err(self.cut(fields)),
        }
    }

    /// The error of the first of `fields` (name and bytes, from here on) the payload cuts.
    #[cold]
    #[inline(never)]
    fn cut(&self, fields: &[(&'static str, usize)]) -> UbxError {
        let mut offset = self.pos;
        for &(field, width) in fields {
            if offset + width > self.payload.len() {
                let detail = Detail::Short { offset, width, length: self.payload.len() };
                return self.error(UbxErrorKind::ShortPayload, field, detail);
            }
            offset += width;
        }
        let (field, width) = fields.last().copied().unwrap_or(("", 0));
        let detail = Detail::Short { offset: offset - width, width, length: self.payload.len() };
        self.error(UbxErrorKind::ShortPayload, field, detail)
    }

    /// The bytes left after `after` bytes the layout still takes (a field of the bytes left).
    pub fn left(&mut self, after: usize) -> &'a [u8] {
        let width = self.remaining().saturating_sub(after);
        let bytes = &self.payload[self.pos..self.pos + width];
        self.pos += width;
        bytes
    }

    /// The bytes after the layout, as sent.
    pub fn rest(&mut self) -> &'a [u8] {
        self.left(0)
    }

    /// A group's entries: `count` of them (None: as many as the bytes left before `after` bytes
    /// hold, at most `max`), at least `min`.
    pub fn group<E: Entry<'a>>(
        &mut self,
        count: Option<usize>,
        min: usize,
        max: usize,
        after: usize,
        field: &'static str,
    ) -> Result<Group<'a, E>, UbxError> {
        let left = self.remaining();
        let at_least = count.is_none();
        let count = count.unwrap_or_else(|| max.min(left.saturating_sub(after) / E::WIDTH));
        if count < min || count * E::WIDTH > left {
            // A count from the bytes left says the least a group takes (as Python says it).
            let count = if at_least { min } else { count };
            return Err(self.error(
                UbxErrorKind::ShortPayload,
                field,
                Detail::FewEntries { count, at_least, width: E::WIDTH, left },
            ));
        }
        let bytes = self.bytes(count * E::WIDTH, field)?;
        Ok(Group { bytes, stride: 0, entry: PhantomData })
    }

    /// A group's entries of `stride` bytes each (SBF's SBLength: at least the entry's fields,
    /// whose last, its trailing bytes, takes the rest; the field `stride_field` holds it): `count` of
    /// them (None: as many as the bytes left before `after` bytes hold, at most `max`), at least `min`.
    #[allow(clippy::too_many_arguments)]
    pub fn group_strided<E: Entry<'a>>(
        &mut self,
        count: Option<usize>,
        stride: usize,
        min: usize,
        max: usize,
        after: usize,
        field: &'static str,
        stride_field: &'static str,
    ) -> Result<Group<'a, E>, UbxError> {
        if count != Some(0) && stride < E::WIDTH {
            // (the stride of no entry says nothing)
            let detail = Detail::Stride { stride, group: field, width: E::WIDTH };
            return Err(self.error(UbxErrorKind::BadValue, stride_field, detail));
        }
        let left = self.remaining();
        let at_least = count.is_none();
        let count = count.unwrap_or_else(|| max.min(left.saturating_sub(after) / stride));
        if count < min || count * stride > left {
            let count = if at_least { min } else { count };
            return Err(self.error(
                UbxErrorKind::ShortPayload,
                field,
                Detail::FewEntries { count, at_least, width: stride, left },
            ));
        }
        let bytes = self.bytes(count * stride, field)?;
        Ok(Group { bytes, stride, entry: PhantomData })
    }

    /// A group's `count` entries of `stride` bytes (the field `stride_field`), each followed by the
    /// entries of its own group (`nested`, counted by a field of the entry, `inner` bytes each: the
    /// field `inner_field`): SBF's Type-1 sub-blocks and their Type-2. Checked entry by entry, as
    /// Python reads them: a stride shorter than the fields, a count that runs past the payload.
    #[allow(clippy::too_many_arguments)]
    pub fn group_nesting<E: Entry<'a>>(
        &mut self,
        count: usize,
        stride: usize,
        inner: usize,
        field: &'static str,
        stride_field: &'static str,
        nested: &'static str,
        inner_field: &'static str,
    ) -> Result<Nesting<'a, E>, UbxError> {
        if count != 0 && stride < E::WIDTH {
            let detail = Detail::Stride { stride, group: field, width: E::WIDTH };
            return Err(self.error(UbxErrorKind::BadValue, stride_field, detail));
        }
        let left = self.remaining();
        if count * stride > left {
            let detail = Detail::FewEntries { count, at_least: false, width: stride, left };
            return Err(self.error(UbxErrorKind::ShortPayload, field, detail));
        }
        let mut at = 0;
        for k in 0..count {
            let rest = left - at;
            if stride > rest {
                let detail = Detail::FewEntries { count: count - k, at_least: false, width: stride, left: rest };
                return Err(self.error(UbxErrorKind::ShortPayload, field, detail));
            }
            let n = E::nested_count(&self.payload[self.pos + at..self.pos + at + stride]);
            at += stride;
            if n != 0 && inner < E::NESTED_WIDTH {
                let detail = Detail::Stride { stride: inner, group: nested, width: E::NESTED_WIDTH };
                return Err(self.error(UbxErrorKind::BadValue, inner_field, detail));
            }
            if n * inner > left - at {
                let detail = Detail::FewEntries { count: n, at_least: false, width: inner, left: left - at };
                return Err(self.error(UbxErrorKind::ShortPayload, nested, detail));
            }
            at += n * inner;
        }
        let bytes = self.bytes(at, field)?;
        Ok(Nesting { bytes, count, stride, inner, entry: PhantomData })
    }
}

/// A payload being written into a caller's buffer, little endian.
#[derive(Debug)]
pub struct ByteWriter<'b> {
    buf: &'b mut [u8],
    len: usize,
    overflow: usize,
    protocol: &'static str,
}

impl<'b> ByteWriter<'b> {
    /// A writer at the start of `buf`.
    pub fn new(buf: &'b mut [u8]) -> Self {
        ByteWriter { buf, len: 0, overflow: 0, protocol: "UBX" }
    }

    /// The bytes written (or that would have been, past the buffer's end).
    pub fn len(&self) -> usize {
        self.len + self.overflow
    }

    /// Whether nothing was written.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Writes `bytes` (past the buffer's end, counts them only: `len` says what it takes).
    pub fn put(&mut self, bytes: &[u8]) {
        match self.buf.get_mut(self.len..self.len + bytes.len()) {
            Some(slot) if self.overflow == 0 => {
                slot.copy_from_slice(bytes);
                self.len += bytes.len();
            }
            _ => self.overflow += bytes.len(),
        }
    }

    /// Writes the characters or bytes of a field of `width` bytes (None: any).
    pub fn put_sized(
        &mut self,
        bytes: &[u8],
        width: Option<usize>,
        message: &'static str,
        field: &'static str,
    ) -> Result<(), UbxError> {
        match width {
            Some(expected) if expected != bytes.len() => Err(UbxError {
                kind: UbxErrorKind::BadValue,
                protocol: self.protocol,
                message,
                class_id: None,
                field: Some(field),
                detail: Detail::Size { expected, found: bytes.len() },
            }),
            _ => {
                self.put(bytes);
                Ok(())
            }
        }
    }
}

/// Writes the frame of class `class`, id `id` whose payload `payload` writes, into `buf`: sync,
/// class, id, length, payload and checksum; the frame's bytes.
pub fn encode_frame<'b>(
    buf: &'b mut [u8],
    class: u8,
    id: u8,
    message: &'static str,
    payload: impl FnOnce(&mut ByteWriter<'_>) -> Result<(), UbxError>,
) -> Result<&'b [u8], UbxError> {
    let room = buf.len().saturating_sub(HEADER_SIZE + CHECKSUM_SIZE);
    let (head, body) = buf.split_at_mut(buf.len().min(HEADER_SIZE));
    let mut w = ByteWriter::new(&mut body[..room]);
    payload(&mut w)?;
    let length = w.len();
    let need = HEADER_SIZE + length + CHECKSUM_SIZE;
    if length > MAX_PAYLOAD || w.overflow > 0 || head.len() < HEADER_SIZE {
        return Err(UbxError {
            kind: UbxErrorKind::BufferTooSmall,
            protocol: "UBX",
            message,
            class_id: Some((class, id)),
            field: None,
            detail: Detail::Buffer { need, have: buf.len() },
        });
    }
    let [low, high] = (length as u16).to_le_bytes();
    buf[..HEADER_SIZE].copy_from_slice(&[SYNC[0], SYNC[1], class, id, low, high]);
    let sum = fletcher8(&buf[2..HEADER_SIZE + length]);
    buf[HEADER_SIZE + length..need].copy_from_slice(&sum);
    Ok(&buf[..need])
}

/// Whether a protocol's frames carry the message's key in their header (CASIC's class and id)
/// rather than as the payload's first bytes (SkyTraq's and SiRF's id).
pub fn key_in_header(f: &FrameFormat) -> bool {
    f.identity.iter().all(|&(_, at, bits)| (at + bits).div_ceil(8) <= f.header)
}

/// The protocol's name in errors: `SKYTRAQ`.
fn upper(f: &FrameFormat) -> &'static str {
    match f.name {
        "skytraq" => "SKYTRAQ",
        "sirf" => "SIRF",
        "casic" => "CASIC",
        "rtcm3" => "RTCM3",
        _ => "UBX",
    }
}

/// The header (sync bytes to the payload) and payload of one whole frame of `protocol` (SkyTraq,
/// SiRF, CASIC: the framing of spec/binary/<protocol>/protocol.yaml), its sync bytes, length,
/// checksum and end bytes checked (the Python runtime's `binary.decode_frame`).
pub fn split_frame_of(protocol: Protocol, data: &[u8]) -> Result<(&[u8], &[u8]), UbxError> {
    let f = protocol.framing();
    let name = upper(f);
    let error = |kind, detail| UbxError { kind, protocol: name, message: "", class_id: None, field: None, detail };
    let sync = data.len().min(f.sync_len);
    if data[..sync] != f.sync[..sync] {
        let mut sent = [0u8; 3];
        sent[..sync].copy_from_slice(&data[..sync]);
        let (expected, want) = (f.sync, f.sync_len);
        return Err(error(UbxErrorKind::BadSync, Detail::Sync { expected, want, sent, len: sync }));
    }
    if data.len() < f.header {
        return Err(error(UbxErrorKind::ShortFrame, Detail::Header { need: f.header, have: data.len() }));
    }
    let size = f.frame_len(data);
    let detail = Detail::Length { size, have: data.len() };
    if data.len() != size {
        let kind = if data.len() < size { UbxErrorKind::ShortFrame } else { UbxErrorKind::LongFrame };
        return Err(error(kind, detail));
    }
    let body = size - f.trailer_len();
    let (sent, computed) = f.check(data);
    if sent != computed {
        return Err(error(UbxErrorKind::BadChecksum, Detail::CheckEnd { sent, computed, width: f.trailer_len() }));
    }
    Ok((&data[..f.header], &data[f.header..body]))
}

/// The members of an unknown message's key, the header's bytes `key` (CASIC's class and id, SBF's
/// id): each identity field of the protocol's framing by its name (`class`, `id`; `number`,
/// `revision`), its bits read in the protocol's byte order.
pub fn json_key<W: Write>(j: &mut JsonObject<'_, W>, protocol: Protocol, key: &[u8]) -> fmt::Result {
    let f = protocol.framing();
    let first = f.identity.iter().map(|&(_, at, _)| at).min().unwrap_or(0) / 8;
    let word = |be: bool| {
        key.iter()
            .enumerate()
            .fold(0u32, |w, (i, &b)| if be { w << 8 | u32::from(b) } else { w | u32::from(b) << (8 * i) })
    };
    for &(name, at, bits) in f.identity {
        if (at + bits).div_ceil(8) - first > key.len() {
            continue;
        }
        let shift = if f.big_endian { 8 * key.len() - (at - 8 * first) - bits } else { at - 8 * first };
        j.int(name, (word(f.big_endian) >> shift) & ((1u32 << bits) - 1))?;
    }
    Ok(())
}

/// Writes the frame of `protocol` (SkyTraq, SiRF, CASIC, SBF) of the message told by `key` (class
/// and id in CASIC's header, the id in SBF's; the id, and sub-id, before the fields in SkyTraq's
/// and SiRF's payload)
/// whose fields `payload` writes, into `buf`: sync, header, payload, checksum and end bytes.
pub fn encode_frame_of<'b>(
    buf: &'b mut [u8],
    protocol: Protocol,
    key: &[u8],
    message: &'static str,
    payload: impl FnOnce(&mut ByteWriter<'_>) -> Result<(), UbxError>,
) -> Result<&'b [u8], UbxError> {
    encode_frame_with(buf, protocol, key, message, |_| {}, payload)
}

/// [`encode_frame_of`] with the header's other fields (Unicore's time and status, which a decoded
/// message keeps): `header` sets them in the frame's header (sync bytes to the payload, zeros but
/// for the sync, length and key) before the checksum is computed.
pub fn encode_frame_with<'b>(
    buf: &'b mut [u8],
    protocol: Protocol,
    key: &[u8],
    message: &'static str,
    header: impl FnOnce(&mut [u8]),
    payload: impl FnOnce(&mut ByteWriter<'_>) -> Result<(), UbxError>,
) -> Result<&'b [u8], UbxError> {
    let f = protocol.framing();
    let in_header = key_in_header(f);
    let room = buf.len().saturating_sub(f.header + f.trailer_len());
    let (head, body) = buf.split_at_mut(buf.len().min(f.header));
    let mut w = ByteWriter { protocol: upper(f), ..ByteWriter::new(&mut body[..room]) };
    if !in_header {
        w.put(key);
    }
    payload(&mut w)?;
    let need = f.header + w.len() + f.trailer_len();
    let length = need - f.length_adds; // the payload's bytes, or the whole frame's (SBF)
    if length > usize::from(f.length_mask) || w.overflow > 0 || head.len() < f.header {
        return Err(UbxError {
            kind: UbxErrorKind::BufferTooSmall,
            protocol: upper(f),
            message,
            class_id: None,
            field: None,
            detail: Detail::Buffer { need, have: buf.len() },
        });
    }
    buf[..f.header].fill(0);
    buf[..f.sync_len].copy_from_slice(&f.sync[..f.sync_len]);
    let field = &mut buf[f.length_at..f.length_at + f.length_size];
    let length = length as u16;
    match (f.length_size, f.big_endian) {
        (2, true) => field.copy_from_slice(&length.to_be_bytes()),
        (2, false) => field.copy_from_slice(&length.to_le_bytes()),
        _ => field[0] = length as u8,
    }
    if in_header {
        // the header's bytes of the key (class and id; SBF: the id of its block number and revision)
        let at = f.identity.iter().map(|&(_, at, _)| at / 8).min().unwrap_or(f.header);
        buf[at..at + key.len()].copy_from_slice(key);
    }
    header(&mut buf[..f.header]);
    let body = need - f.trailer_len();
    let (_, check) = f.check(&buf[..need]); // the checksum of what it covers, and the end bytes
    let (at, end) = if f.check_at == 0 {
        (body, need) // checksum and end bytes after the payload
    } else {
        buf[body..need].copy_from_slice(f.end);
        (f.check_at, f.check_at + f.check_size) // the checksum in the header (SBF)
    };
    let check = if f.check_at == 0 { check } else { check >> (8 * f.end.len()) };
    for (i, slot) in buf[at..end].iter_mut().rev().enumerate() {
        *slot = (check >> (8 * i)) as u8;
    }
    Ok(&buf[..need])
}

/// One entry of a repeated group (a struct generated from the spec): its fixed width, read from
/// and written to exactly that many bytes.
pub trait Entry<'a>: Sized {
    /// The entry's bytes.
    const WIDTH: usize;
    /// The entry of `bytes` (`WIDTH` of them).
    fn read(r: &mut ByteReader<'a>) -> Result<Self, UbxError>;
    /// Writes the entry's fields.
    fn write(&self, w: &mut ByteWriter<'_>) -> Result<(), UbxError>;
    /// The members of its decoded JSON, in order.
    fn json_members<W: Write>(&self, j: &mut JsonObject<'_, W>) -> fmt::Result;
    /// An entry that ends with a group of its own (SBF's Type-2 sub-blocks after a Type-1, a
    /// [`Nesting`]'s): that group's number of entries, from the entry's fields' bytes (`head`, at
    /// least `WIDTH`); 0 for the others.
    fn nested_count(_head: &[u8]) -> usize {
        0
    }
    /// The least bytes of an entry of the group it ends with (0: it ends with none).
    const NESTED_WIDTH: usize = 0;
    /// Sets the group it ends with to the entries of `bytes`, `stride` bytes each (none for
    /// an entry that ends with no group).
    fn set_nested(&mut self, _bytes: &'a [u8], _stride: usize) {}
}

/// The entries of a repeated group, as sent: a view of their bytes, each entry read when asked
/// (from its `stride` bytes: 0 for the entry's width; SBF's SBLength, the entry's fields then its
/// trailing bytes).
pub struct Group<'a, E> {
    bytes: &'a [u8],
    stride: usize,
    entry: PhantomData<E>,
}

/// Entries as the JSON array member `name` of `j`, each an object of its members.
fn json_entries<'a, W: Write, E: Entry<'a>>(
    j: &mut JsonObject<'_, W>,
    name: &str,
    entries: impl Iterator<Item = E>,
) -> fmt::Result {
    let out = j.key(name)?;
    out.write_char('[')?;
    for (i, entry) in entries.enumerate() {
        if i > 0 {
            out.write_char(',')?;
        }
        let mut e = JsonObject::new(&mut *out)?;
        entry.json_members(&mut e)?;
        e.finish()?;
    }
    out.write_char(']')
}

impl<'a, E: Entry<'a>> Group<'a, E> {
    /// The entries of `bytes`, whole entries only (None for a length that is not a whole
    /// number of entries).
    pub fn new(bytes: &'a [u8]) -> Option<Self> {
        (bytes.len().checked_rem(E::WIDTH) == Some(0)).then_some(Group { bytes, stride: 0, entry: PhantomData })
    }

    /// The entries of `bytes`, `stride` bytes each, at least an entry's fields (None for a stride
    /// shorter, or a length that is not a whole number of entries).
    pub fn with_stride(bytes: &'a [u8], stride: usize) -> Option<Self> {
        (stride >= E::WIDTH.max(1) && bytes.len().checked_rem(stride) == Some(0)).then_some(Group {
            bytes,
            stride,
            entry: PhantomData,
        })
    }

    /// The bytes of an entry.
    pub fn stride(&self) -> usize {
        if self.stride == 0 {
            E::WIDTH.max(1)
        } else {
            self.stride
        }
    }

    /// The number of entries.
    pub fn len(&self) -> usize {
        self.bytes.len() / self.stride()
    }

    /// Whether there is none.
    pub fn is_empty(&self) -> bool {
        self.bytes.is_empty()
    }

    /// The entries' bytes, as sent.
    pub fn bytes(&self) -> &'a [u8] {
        self.bytes
    }

    /// The entry at `index`.
    pub fn get(&self, index: usize) -> Option<E> {
        let stride = self.stride();
        let bytes = self.bytes.get(index * stride..(index + 1) * stride)?;
        E::read(&mut ByteReader::new(bytes, "", (0, 0))).ok()
    }

    /// The entries, in order.
    pub fn iter(&self) -> impl Iterator<Item = E> + 'a {
        self.bytes.chunks_exact(self.stride()).filter_map(|bytes| E::read(&mut ByteReader::new(bytes, "", (0, 0))).ok())
    }

    /// Writes the entries.
    pub fn write(&self, w: &mut ByteWriter<'_>) {
        w.put(self.bytes);
    }

    /// Writes the entries of a stride whose field (`stride_field`) says `stride` bytes: an error
    /// when the entries are of another size.
    pub fn write_strided(
        &self,
        w: &mut ByteWriter<'_>,
        stride: usize,
        message: &'static str,
        stride_field: &'static str,
        field: &'static str,
    ) -> Result<(), UbxError> {
        if !self.is_empty() && self.stride() != stride {
            return Err(UbxError {
                kind: UbxErrorKind::BadValue,
                protocol: w.protocol,
                message,
                class_id: None,
                field: Some(stride_field),
                detail: Detail::StrideWritten { written: self.stride(), group: field, stride },
            });
        }
        w.put(self.bytes);
        Ok(())
    }

    /// The entries as a JSON array member.
    pub fn json<W: Write>(&self, j: &mut JsonObject<'_, W>, name: &str) -> fmt::Result {
        json_entries(j, name, self.iter())
    }
}

impl<E> Clone for Group<'_, E> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<E> Copy for Group<'_, E> {}

impl<E> Default for Group<'_, E> {
    fn default() -> Self {
        Group { bytes: &[], stride: 0, entry: PhantomData }
    }
}

impl<E> PartialEq for Group<'_, E> {
    fn eq(&self, other: &Self) -> bool {
        self.bytes == other.bytes && self.stride == other.stride
    }
}

impl<'a, E: Entry<'a> + fmt::Debug> fmt::Debug for Group<'a, E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

/// The entries of a group whose entries each end with a group of their own (SBF's Type-1
/// sub-blocks of SB1Length, each followed by its N2 Type-2 sub-blocks of SB2Length), as sent: a view
/// of their bytes, each entry (and its own group, a [`Group`] of `inner`-byte entries) read when
/// asked, nothing allocated.
pub struct Nesting<'a, E> {
    bytes: &'a [u8],
    count: usize,
    stride: usize,
    inner: usize,
    entry: PhantomData<E>,
}

impl<'a, E: Entry<'a>> Nesting<'a, E> {
    /// The `count` entries of `bytes`: each `stride` bytes (at least its fields'), then its own
    /// group's entries of `inner` bytes each (None when `bytes` is not exactly that).
    pub fn new(bytes: &'a [u8], count: usize, stride: usize, inner: usize) -> Option<Self> {
        let mut at = 0;
        for _ in 0..count {
            let head = bytes.get(at..at + stride).filter(|_| stride >= E::WIDTH.max(1))?;
            let n = E::nested_count(head);
            if n != 0 && inner < E::NESTED_WIDTH.max(1) {
                return None;
            }
            at += stride + n * inner;
        }
        (at == bytes.len()).then_some(Nesting { bytes, count, stride, inner, entry: PhantomData })
    }

    /// The number of entries.
    pub fn len(&self) -> usize {
        self.count
    }

    /// Whether there is none.
    pub fn is_empty(&self) -> bool {
        self.count == 0
    }

    /// The bytes of every entry and of their groups' entries, as sent.
    pub fn bytes(&self) -> &'a [u8] {
        self.bytes
    }

    /// The bytes of an entry (its fields, then its trailing bytes), of an entry of an entry's group.
    pub fn strides(&self) -> (usize, usize) {
        (self.stride, self.inner)
    }

    /// The entries, in order (each with its own group's).
    pub fn iter(&self) -> impl Iterator<Item = E> + 'a {
        let (bytes, stride, inner) = (self.bytes, self.stride, self.inner);
        let mut at = 0;
        (0..self.count).map_while(move |_| {
            let head = bytes.get(at..at + stride)?;
            let end = at + stride + E::nested_count(head) * inner;
            let mut entry = E::read(&mut ByteReader::new(head, "", (0, 0))).ok()?;
            entry.set_nested(bytes.get(at + stride..end)?, inner);
            at = end;
            Some(entry)
        })
    }

    /// The entry at `index` (its entries before it are walked over).
    pub fn get(&self, index: usize) -> Option<E> {
        self.iter().nth(index)
    }

    /// Whether an entry's own group has entries.
    fn has_inner(&self) -> bool {
        let mut at = 0;
        for _ in 0..self.count {
            let Some(head) = self.bytes.get(at..at + self.stride) else { return false };
            let n = E::nested_count(head);
            if n != 0 {
                return true;
            }
            at += self.stride;
        }
        false
    }

    /// Writes the entries when they are of the strides the message's fields say (`stride_field`
    /// `stride` for those of `field`, `inner_field` `inner` for those of their groups, `nested`);
    /// an error naming the field they differ from otherwise.
    #[allow(clippy::too_many_arguments)]
    pub fn write_strided(
        &self,
        w: &mut ByteWriter<'_>,
        (stride, inner): (usize, usize),
        message: &'static str,
        (stride_field, inner_field): (&'static str, &'static str),
        field: &'static str,
        nested: &'static str,
    ) -> Result<(), UbxError> {
        let wrong = if !self.is_empty() && self.stride != stride {
            Some((stride_field, field, self.stride, stride))
        } else if self.inner != inner && self.has_inner() {
            Some((inner_field, nested, self.inner, inner))
        } else {
            None
        };
        if let Some((name, group, written, stride)) = wrong {
            return Err(UbxError {
                kind: UbxErrorKind::BadValue,
                protocol: w.protocol,
                message,
                class_id: None,
                field: Some(name),
                detail: Detail::StrideWritten { written, group, stride },
            });
        }
        w.put(self.bytes);
        Ok(())
    }

    /// The entries as a JSON array member (each entry's members, its own group's last).
    pub fn json<W: Write>(&self, j: &mut JsonObject<'_, W>, name: &str) -> fmt::Result {
        json_entries(j, name, self.iter())
    }
}

impl<E> Clone for Nesting<'_, E> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<E> Copy for Nesting<'_, E> {}

impl<E> Default for Nesting<'_, E> {
    fn default() -> Self {
        Nesting { bytes: &[], count: 0, stride: 0, inner: 0, entry: PhantomData }
    }
}

impl<E> PartialEq for Nesting<'_, E> {
    fn eq(&self, other: &Self) -> bool {
        (self.bytes, self.count, self.stride, self.inner) == (other.bytes, other.count, other.stride, other.inner)
    }
}

impl<'a, E: Entry<'a> + fmt::Debug> fmt::Debug for Nesting<'a, E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

/// A float field with special values (SBF's do-not-use -2e10): its value, or the special value whose
/// bit pattern (in the field's own width, widened) it holds; `specials` are (bits, id).
pub fn float_reading(bits: u64, value: f64, specials: &[(u64, &'static str)]) -> super::ais::Reading<f64> {
    specials
        .iter()
        .find(|&&(raw, _)| raw == bits)
        .map_or(super::ais::Reading::Value(value), |&(_, id)| super::ais::Reading::Special(id))
}

/// A float member: a double as Python's `repr` writes it ([`write_repr`](super::repr::write_repr)), NaN
/// and the infinities as the strings `"nan"`, `"inf"`, `"-inf"`.
pub fn json_float<W: Write>(j: &mut JsonObject<'_, W>, name: &str, value: f64) -> fmt::Result {
    let out = j.key(name)?;
    if value.is_nan() {
        return out.write_str("\"nan\"");
    }
    if value.is_infinite() {
        return out.write_str(if value > 0.0 { "\"inf\"" } else { "\"-inf\"" });
    }
    super::repr::write_repr(out, value)
}

/// A characters member: the bytes as ISO 8859-1 text, escaped as Python's `json.dumps` escapes
/// (ensure_ascii: `\n`, `\r`, `\t`, `\b`, `\f`, and `\u00hh` outside 0x20-0x7E).
pub fn json_chars<W: Write>(j: &mut JsonObject<'_, W>, name: &str, value: &[u8]) -> fmt::Result {
    let out = j.key(name)?;
    out.write_char('"')?;
    for &byte in value {
        match byte {
            b'"' => out.write_str("\\\"")?,
            b'\\' => out.write_str("\\\\")?,
            b'\n' => out.write_str("\\n")?,
            b'\r' => out.write_str("\\r")?,
            b'\t' => out.write_str("\\t")?,
            0x08 => out.write_str("\\b")?,
            0x0C => out.write_str("\\f")?,
            0x20..=0x7E => out.write_char(char::from(byte))?,
            _ => write!(out, "\\u{:04x}", byte)?,
        }
    }
    out.write_char('"')
}

/// A bytes member: lower-case hex.
pub fn json_hex<W: Write>(j: &mut JsonObject<'_, W>, name: &str, value: &[u8]) -> fmt::Result {
    let out = j.key(name)?;
    out.write_char('"')?;
    value.iter().try_for_each(|byte| write!(out, "{byte:02x}"))?;
    out.write_char('"')
}

#[cfg(test)]
mod tests {
    use super::*;
    extern crate std;
    use std::string::{String, ToString};

    const ACK: [u8; 10] = [0xB5, 0x62, 0x05, 0x01, 0x02, 0x00, 0x06, 0x00, 0x0E, 0x37];

    #[test]
    fn a_frame_splits_into_class_id_and_payload() {
        assert_eq!(split_frame(&ACK), Ok((5, 1, &ACK[6..8])));
        assert_eq!(fletcher8(&ACK[2..8]), [0x0E, 0x37]);
    }

    #[test]
    fn fletcher8_eight_bytes_a_step_sums_as_byte_by_byte() {
        let data: std::vec::Vec<u8> = (0u32..700).map(|i| (i.wrapping_mul(2_654_435_761) >> 13) as u8 | 0x80).collect();
        for end in 0..data.len() {
            for start in [0, 1, 7] {
                let (mut a, mut b) = (0u8, 0u8);
                for &byte in &data[start.min(end)..end] {
                    a = a.wrapping_add(byte);
                    b = b.wrapping_add(a);
                }
                assert_eq!(fletcher8(&data[start.min(end)..end]), [a, b], "bytes {start}..{end}");
            }
        }
        assert_eq!(fletcher8(&[0xFF; 300]), [0xD4, 0xA2]);
    }

    #[test]
    fn frame_errors_say_what_is_wrong() {
        let mut bad = ACK;
        bad[9] = 0x38;
        let err = split_frame(&bad).unwrap_err();
        assert_eq!(err.to_string(), "bad_checksum: UBX 0x05 0x01: checksum 0E 38, computed 0E 37");
        let err = split_frame(&ACK[..9]).unwrap_err();
        assert_eq!(err.to_string(), "short_frame: UBX 0x05 0x01: the length field says 10 bytes, the frame has 9");
        assert_eq!(
            split_frame(&[0xB5, 0x00]).unwrap_err().text().to_string(),
            "a UBX frame starts with B5 62, not B5 00"
        );
        assert_eq!(split_frame(&ACK[..4]).unwrap_err().kind, UbxErrorKind::ShortFrame);
    }

    #[test]
    fn a_run_of_fields_checks_its_length_once_and_names_the_field_cut() {
        let fields = [("itow", 4), ("year", 2), ("month", 1)];
        let mut r = ByteReader::new(&[1, 0, 0, 0, 0xEA, 7, 3, 9], "NAV-PVT", (1, 7));
        assert_eq!(r.run::<7>(&fields), Ok(&[1, 0, 0, 0, 0xEA, 7, 3]));
        assert_eq!(r.remaining(), 1);
        for (length, field, text) in [
            (0, "itow", "itow needs bytes 0-3, the payload has 0"),
            (5, "year", "year needs bytes 4-5, the payload has 5"),
            (6, "month", "month needs byte 6, the payload has 6"),
        ] {
            let payload = [0u8; 7];
            let err = ByteReader::new(&payload[..length], "NAV-PVT", (1, 7)).run::<7>(&fields).unwrap_err();
            assert_eq!((err.kind, err.field), (UbxErrorKind::ShortPayload, Some(field)));
            assert_eq!(err.text().to_string(), text);
        }
    }

    #[test]
    fn a_short_payload_names_field_and_bytes() {
        let mut r = ByteReader::new(&[0; 28], "NAV-PVT", (1, 7));
        r.bytes(28, "head").unwrap();
        let err = r.array::<4>("lat").unwrap_err();
        assert_eq!(err.to_string(), "short_payload: UBX NAV-PVT: lat needs bytes 28-31, the payload has 28");
    }

    #[test]
    fn a_frame_is_written_with_length_and_checksum() {
        let mut buf = [0u8; 16];
        let frame = encode_frame(&mut buf, 5, 1, "ACK-ACK", |w| {
            w.put(&[6, 0]);
            Ok(())
        });
        assert_eq!(frame, Ok(&ACK[..]));
        let mut small = [0u8; 9];
        let err = encode_frame(&mut small, 5, 1, "ACK-ACK", |w| {
            w.put(&[6, 0]);
            Ok(())
        });
        assert_eq!(err.unwrap_err().kind, UbxErrorKind::BufferTooSmall);
    }

    #[test]
    fn floats_are_written_as_python_writes_them() {
        let cases = [
            (0.0, "0.0"),
            (1e-5, "1e-05"),
            (1.5e16, "1.5e+16"),
            (0.25, "0.25"),
            (f64::NAN, "\"nan\""),
            (-0.0, "-0.0"),
            (100.0, "100.0"),
            (1234567890123456.0, "1234567890123456.0"),
            (0.000123, "0.000123"),
            (-2.5e-300, "-2.5e-300"),
            (1e22, "1e+22"),
            // A float widened to a double, halfway between two 17-digit decimals: ties to even.
            (f64::from(3.912_788_4_f32), "3.9127883911132812"),
        ];
        for (value, text) in cases {
            let mut out = String::new();
            let mut j = JsonObject::new(&mut out).unwrap();
            json_float(&mut j, "x", value).unwrap();
            j.finish().unwrap();
            assert_eq!(out, std::format!("{{\"x\":{text}}}"));
        }
    }
}
