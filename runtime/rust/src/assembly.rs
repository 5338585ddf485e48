//! AIS messages assembled across sentences, as Python's `nmeaspec.assembly` assembles them (the
//! shared cases are tests/data/ais/assembly_cases.jsonl), in fixed memory: `SLOTS` messages under
//! way at once, each holding up to `CAPACITY` bytes of payload.
//!
//! A message of one sentence comes back at once. A message of several comes back with its last
//! missing fragment, in whatever order they came, interleaved with any other sentences; it is
//! joined under its key: the TAG group (with its source) when the line has one, else the talker,
//! sentence, channel and sequential message id. A message that cannot complete is given up as
//! incomplete with the fragments that came: when a fragment it has comes again or one with
//! another count, when `lifetime` more encapsulation sentences have come since its first
//! fragment, when every slot is taken and a newer message needs one (the oldest goes), when its
//! payload outgrows `CAPACITY` or its key [`KEY_CAPACITY`], and at [`Assembler::finish`].
//!
//! Each message names its sentences by the indices of the lines fed ([`Assembler::feed`] counts
//! every line from 0), in fragment order, so that the caller writes back exactly what came.

use core::fmt;

use super::{Number, Sign, TagBlocks};

/// The most fragments of one message (NMEA 0183: a count is one digit).
pub const MAX_FRAGMENTS: usize = 9;
/// The bytes of a key: a TAG source and group id, or a talker, sentence, channel and id.
pub const KEY_CAPACITY: usize = 40;

/// What an encapsulation sentence (`!AIVDM`) says of the message it carries all or part of: the
/// fields its spec's `encapsulates` names, with its talker and sentence for the key.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Fragment<'a> {
    /// The talker (`AI`) and the sentence id (`VDM`), for the key.
    pub talker: &'a str,
    #[allow(missing_docs)]
    pub sentence: &'a str,
    /// How many fragments the message has (1 to [`MAX_FRAGMENTS`]), and which this is.
    pub count: u8,
    #[allow(missing_docs)]
    pub number: u8,
    /// The sequential message id and the radio channel, for the key.
    pub sequence: Option<u8>,
    #[allow(missing_docs)]
    pub channel: Option<&'a str>,
    /// The armored payload (of this fragment) and its fill bits.
    pub payload: &'a str,
    #[allow(missing_docs)]
    pub fill_bits: u8,
}

impl<'a> Fragment<'a> {
    /// From an encapsulation sentence's talker and sentence id, its count, number, sequential id
    /// and fill bits, channel and payload; `None` when the count is not 1 to [`MAX_FRAGMENTS`] or
    /// the number is empty. A number counts when it is a whole 0-255 written without a minus: the
    /// sequential id is `None` otherwise, the fill bits 0.
    pub fn of(
        (talker, sentence): (&'a str, &'a str),
        [count, number, sequence, fill_bits]: [Option<Number>; 4],
        channel: Option<&'a str>,
        payload: Option<&'a str>,
    ) -> Option<Self> {
        // a whole 0-255 written without a minus
        let small = |n: Number| u8::try_from(n.digits).ok().filter(|_| n.scale == 0 && n.sign != Sign::Minus);
        let count = small(count?).filter(|c| (1..=MAX_FRAGMENTS as u8).contains(c))?;
        Some(Self {
            talker,
            sentence,
            count,
            number: small(number?)?,
            sequence: sequence.and_then(small),
            channel,
            payload: payload.unwrap_or_default(),
            fill_bits: fill_bits.and_then(small).unwrap_or_default(),
        })
    }
}

/// A message done with: the lines that carried it and, when it is whole, its payload and fill
/// bits (`None`: given up as incomplete, `incomplete_message`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Assembled<'e> {
    /// The indices of the lines fed that carried it, in fragment order.
    pub lines: &'e [u32],
    /// Their fragment numbers, and how many fragments the message has.
    pub numbers: &'e [u8],
    #[allow(missing_docs)]
    pub count: u8,
    /// The joined payload and the last fragment's fill bits.
    pub joined: Option<(&'e str, u8)>,
}

impl Assembled<'_> {
    /// The message of a given-up message's `incomplete_message` error: `fragment 2 of 2 never
    /// came`, `fragments 1, 3 of 3 never came`.
    pub fn incomplete_message(&self) -> impl fmt::Display + '_ {
        Incomplete(self)
    }
}

struct Incomplete<'a, 'e>(&'a Assembled<'e>);

impl fmt::Display for Incomplete<'_, '_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let done = self.0;
        let mut missing = (1..=done.count).filter(|n| !done.numbers.contains(n));
        let several = missing.clone().nth(1).is_some();
        f.write_str(if several { "fragments " } else { "fragment " })?;
        if let Some(first) = missing.next() {
            write!(f, "{first}")?;
        }
        for n in missing {
            write!(f, ", {n}")?;
        }
        write!(f, " of {} never came", done.count)
    }
}

#[derive(Clone, Copy)]
struct Part {
    number: u8,
    line: u32,
    fill_bits: u8,
    start: usize,
    end: usize,
}

const NO_PART: Part = Part { number: 0, line: 0, fill_bits: 0, start: 0, end: 0 };

/// A message under way (`count` 0: a free slot). Payloads are kept in the order they came.
struct Slot<const CAPACITY: usize> {
    key: [u8; KEY_CAPACITY],
    key_len: usize,
    count: u8,
    started: u32,
    parts: [Part; MAX_FRAGMENTS],
    n_parts: usize,
    payload: [u8; CAPACITY],
}

impl<const CAPACITY: usize> Slot<CAPACITY> {
    const FREE: Self = Self {
        key: [0; KEY_CAPACITY],
        key_len: 0,
        count: 0,
        started: 0,
        parts: [NO_PART; MAX_FRAGMENTS],
        n_parts: 0,
        payload: [0; CAPACITY],
    };

    fn key(&self) -> &[u8] {
        &self.key[..self.key_len]
    }

    fn has(&self, number: u8) -> bool {
        self.parts[..self.n_parts].iter().any(|p| p.number == number)
    }

    fn used(&self) -> usize {
        self.parts[..self.n_parts].last().map_or(0, |p| p.end)
    }
}

/// Joins the fragments of multi-sentence AIS messages (see the module's doc).
pub struct Assembler<const SLOTS: usize = 16, const CAPACITY: usize = 558> {
    slots: [Slot<CAPACITY>; SLOTS],
    lifetime: u32,
    lines: u32,
    seen: u32,
    out_lines: [u32; MAX_FRAGMENTS],
    out_numbers: [u8; MAX_FRAGMENTS],
    out_payload: [u8; CAPACITY],
}

impl<const SLOTS: usize, const CAPACITY: usize> Assembler<SLOTS, CAPACITY> {
    /// An assembler that gives a message up when `lifetime` (at least 1) encapsulation sentences
    /// have come since its first fragment.
    pub const fn new(lifetime: u32) -> Self {
        Self {
            slots: [Slot::FREE; SLOTS],
            lifetime,
            lines: 0,
            seen: 0,
            out_lines: [0; MAX_FRAGMENTS],
            out_numbers: [0; MAX_FRAGMENTS],
            out_payload: [0; CAPACITY],
        }
    }

    /// Counts the line and gives `done` what its fragment (`None`: the line carries no AIS
    /// message) completes or gives up, in order; `tags` are the line's TAG blocks.
    pub fn feed(&mut self, fragment: Option<Fragment<'_>>, tags: TagBlocks<'_>, mut done: impl FnMut(Assembled<'_>)) {
        let line = self.lines;
        self.lines = self.lines.wrapping_add(1);
        let Some(fragment) = fragment else { return };
        self.seen = self.seen.wrapping_add(1);
        while let Some(oldest) =
            self.oldest().filter(|&i| self.seen.wrapping_sub(self.slots[i].started) >= self.lifetime)
        {
            self.give_up(oldest, &mut done);
        }
        let (lines, numbers) = ([line], [fragment.number]);
        let alone = |joined| Assembled { lines: &lines, numbers: &numbers, count: fragment.count, joined };
        if fragment.count == 1 {
            return done(alone(Some((fragment.payload, fragment.fill_bits))));
        }
        let mut key = [0; KEY_CAPACITY];
        let Some(key_len) = write_key(&mut key, &fragment, tags) else {
            return done(alone(None));
        };
        let key = &key[..key_len];
        let mut slot = self.slots.iter().position(|s| s.count != 0 && s.key() == key);
        if let Some(i) = slot.filter(|&i| self.slots[i].has(fragment.number) || self.slots[i].count != fragment.count) {
            self.give_up(i, &mut done); // a new message under the same key
            slot = None;
        }
        let i = match slot {
            Some(i) => i,
            None => {
                let free = match self.slots.iter().position(|s| s.count == 0) {
                    Some(free) => free,
                    None => {
                        let Some(oldest) = self.oldest() else {
                            return done(alone(None));
                        };
                        self.give_up(oldest, &mut done);
                        oldest
                    }
                };
                let s = &mut self.slots[free];
                s.key[..key.len()].copy_from_slice(key);
                s.key_len = key.len();
                s.count = fragment.count;
                s.started = self.seen;
                s.n_parts = 0;
                free
            }
        };
        let s = &mut self.slots[i];
        let (start, payload) = (s.used(), fragment.payload.as_bytes());
        if start + payload.len() > CAPACITY {
            if s.n_parts > 0 {
                self.give_up(i, &mut done);
            } else {
                s.count = 0; // a message that never started
            }
            return done(alone(None));
        }
        s.payload[start..start + payload.len()].copy_from_slice(payload);
        s.parts[s.n_parts] =
            Part { number: fragment.number, line, fill_bits: fragment.fill_bits, start, end: start + payload.len() };
        s.n_parts += 1;
        if s.n_parts == usize::from(s.count) {
            let (n, count, used, fill_bits) = self.join(i);
            // Fragments' payloads are text, and joined whole.
            let text = core::str::from_utf8(&self.out_payload[..used]).unwrap_or_default();
            let (lines, numbers) = (&self.out_lines[..n], &self.out_numbers[..n]);
            done(Assembled { lines, numbers, count, joined: Some((text, fill_bits)) });
        }
    }

    /// Gives up every message still under way, oldest first (the stream has ended).
    pub fn finish(&mut self, mut done: impl FnMut(Assembled<'_>)) {
        while let Some(oldest) = self.oldest() {
            self.give_up(oldest, &mut done);
        }
    }

    /// The slot of the message under way that started first.
    fn oldest(&self) -> Option<usize> {
        (0..SLOTS).filter(|&i| self.slots[i].count != 0).min_by_key(|&i| self.slots[i].started)
    }

    fn give_up(&mut self, slot: usize, done: &mut impl FnMut(Assembled<'_>)) {
        let (n, count, _, _) = self.join(slot);
        done(Assembled { lines: &self.out_lines[..n], numbers: &self.out_numbers[..n], count, joined: None });
    }

    /// Frees the slot, its lines, fragment numbers and payload put in fragment order into the
    /// output buffers: how many lines, the fragment count, how many bytes of payload, and the last
    /// fragment's fill bits.
    fn join(&mut self, slot: usize) -> (usize, u8, usize, u8) {
        let s = &mut self.slots[slot];
        let parts = &mut s.parts[..s.n_parts];
        parts.sort_unstable_by_key(|p| p.number);
        let mut used = 0;
        for (k, part) in parts.iter().enumerate() {
            self.out_lines[k] = part.line;
            self.out_numbers[k] = part.number;
            let len = part.end - part.start;
            self.out_payload[used..used + len].copy_from_slice(&s.payload[part.start..part.end]);
            used += len;
        }
        let count = core::mem::take(&mut s.count);
        (s.n_parts, count, used, parts.last().map_or(0, |p| p.fill_bits))
    }
}

/// Writes the fragment's key into `key`: `g`, the TAG source and group id when the line has a
/// group, else `a`, the talker, sentence, channel and sequential id, each ended by a NUL. `None`:
/// it does not fit.
fn write_key(key: &mut [u8; KEY_CAPACITY], fragment: &Fragment<'_>, tags: TagBlocks<'_>) -> Option<usize> {
    let mut len = 0;
    let mut put = |text: &[u8]| -> Option<()> {
        let end = len + text.len() + 1;
        key.get_mut(len..end - 1)?.copy_from_slice(text);
        key[end - 1] = 0;
        len = end;
        Some(())
    };
    if let Some(group) = tags.get("g") {
        // The id is a number (Python compares it as one): leading zeros name the same group.
        let id = group.rsplit('-').next().unwrap_or(group).trim_start_matches('0');
        let id = if id.is_empty() { "0" } else { id };
        put(b"g")?;
        put(tags.get("s").unwrap_or_default().as_bytes())?;
        put(id.as_bytes())?;
    } else {
        put(b"a")?;
        put(fragment.talker.as_bytes())?;
        put(fragment.sentence.as_bytes())?;
        put(fragment.channel.unwrap_or_default().as_bytes())?;
        put(&[u8::from(fragment.sequence.is_some()), fragment.sequence.unwrap_or_default()])?;
    }
    Some(len)
}
