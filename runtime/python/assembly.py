"""AIS messages assembled across sentences.

An AIS message longer than one sentence holds (a type 5 static report, most binary messages)
arrives as fragments: `!AIVDM,2,1,3,B,...,0` then `!AIVDM,2,2,3,B,...,2`, each naming how many
fragments there are, which one it is, a sequential message id (0-9, so that a few messages can be
under way at once) and the radio channel. Behind TAG blocks the fragments may instead be tied
together by a group (`g:1-2-73874`). `MessageAssembler` joins them:

    assembler = MessageAssembler()
    for sentence in nmeaspec.sentences(stream):
        for done in assembler.feed(sentence):
            print(done.message or done.error, [s.to_sentence() for s in done.sentences])
    for done in assembler.finish():     # what was left incomplete when the stream ended
        ...

A message of one sentence comes back at once. A message of several comes back with its last
missing fragment, whatever the order they came in, interleaved with any other sentences; it keeps
its sentences (in fragment order), so it writes back exactly as received. A message that cannot
complete comes back with an `incomplete_message` error and the fragments that came: when a
fragment it has comes again (a new message under its key) or one with another total, when
`lifetime` more encapsulation sentences have come since its first fragment, when every one of
the `slots` is taken and a newer message needs one (the oldest goes), or when its payload would
outgrow `capacity` characters or its key KEY_CAPACITY bytes (the bounds of the C and Rust
assemblers' fixed memory, which give up the same messages). Nothing but the incomplete message is
lost.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, NamedTuple

from .ais import Fragment, Message
from .ais_messages import decode_payload
from .api import Tagged
from .runtime import NmeaError

MAX_FRAGMENTS = 9
"""The most fragments of one message (NMEA 0183: a count is one digit)."""
KEY_CAPACITY = 40
"""The bytes of a key as the C and Rust assemblers keep it (each part ended by a NUL): a TAG
source and group id, or a talker, sentence, channel and sequential id."""


class Assembled(NamedTuple):
    """A message and the sentences that carried it (in fragment order; a Tagged line when it came
    with TAG blocks). `message` is None when `error` says why: the payload did not decode, or the
    message is incomplete (`incomplete_message`)."""

    sentences: tuple[Any, ...]
    message: Message | None
    error: NmeaError | None


@dataclass
class _Partial:
    key: tuple[str, ...]
    total: int
    started: int  # the encapsulation sentence it started with (MessageAssembler's count)
    parts: dict[int, tuple[Any, Fragment]] = field(default_factory=dict)


class MessageAssembler:
    """Joins the fragments of multi-sentence AIS messages (see the module's doc). `slots`: how many
    messages may be under way at once; `lifetime`: how many encapsulation sentences may come after
    a message's first fragment before it is given up."""

    def __init__(self, slots: int = 16, lifetime: int = 100, capacity: int = 558) -> None:
        if slots < 1 or lifetime < 1:
            raise ValueError("slots and lifetime are at least 1")
        self.slots = slots
        self.lifetime = lifetime
        self.capacity = capacity
        self._seen = 0
        self._partials: dict[tuple[str, ...], _Partial] = {}  # in the order they started

    def feed(self, line: Any) -> list[Assembled]:
        """What the sentence (or Tagged line) completes or gives up: nothing for a sentence that
        carries no AIS message, or a fragment of one still under way."""
        sentence = line.sentence if isinstance(line, Tagged) else line
        fragment = getattr(sentence, "fragment", None)
        if fragment is None:
            return []
        self._seen += 1
        done = [self._incomplete(p) for p in list(self._partials.values())
                if self._seen - p.started >= self.lifetime]
        if fragment.total == 1:
            return done + [_decoded((line,), fragment.payload, fragment.fill_bits)]
        key = _key(line, sentence, fragment)
        if key is None:
            return done + [_alone(line, fragment)]
        partial = self._partials.get(key)
        if partial is not None and (fragment.number in partial.parts or fragment.total != partial.total):
            done.append(self._incomplete(partial))  # a new message under the same key
            partial = None
        if partial is None:
            if len(self._partials) >= self.slots:
                done.append(self._incomplete(next(iter(self._partials.values()))))
            partial = self._partials[key] = _Partial(key, fragment.total, self._seen)
        if sum(len(f.payload) for _, f in partial.parts.values()) + len(fragment.payload) > self.capacity:
            if partial.parts:
                done.append(self._incomplete(partial))
            else:
                del self._partials[key]  # a message that never started
            return done + [_alone(line, fragment)]
        partial.parts[fragment.number] = (line, fragment)
        if len(partial.parts) == partial.total:
            del self._partials[key]
            parts = [partial.parts[n] for n in sorted(partial.parts)]
            payload = "".join(f.payload for _, f in parts)
            done.append(_decoded(tuple(s for s, _ in parts), payload, parts[-1][1].fill_bits))
        return done

    def finish(self) -> list[Assembled]:
        """The messages still under way, given up as incomplete (the stream has ended)."""
        return [self._incomplete(p) for p in list(self._partials.values())]

    def _incomplete(self, partial: _Partial) -> Assembled:
        del self._partials[partial.key]
        numbers = sorted(partial.parts)
        return _given_up(tuple(partial.parts[n][0] for n in numbers), numbers, partial.total)


def _given_up(sentences: tuple[Any, ...], numbers: list[int], total: int) -> Assembled:
    missing = [n for n in range(1, total + 1) if n not in numbers]
    error = NmeaError("incomplete_message",
                      f"fragment{'s' * (len(missing) > 1)} {', '.join(map(str, missing))} of {total} never came",
                      "AIS")
    return Assembled(sentences, None, error)


def _alone(line: Any, fragment: Fragment) -> Assembled:
    """A fragment given up on its own: its key or payload does not fit."""
    return _given_up((line,), [fragment.number], fragment.total)


def _decoded(sentences: tuple[Any, ...], payload: str, fill_bits: int) -> Assembled:
    try:
        return Assembled(sentences, decode_payload(payload, fill_bits), None)
    except NmeaError as err:
        return Assembled(sentences, None, err)


def _key(line: Any, sentence: Any, fragment: Fragment) -> tuple[str, ...] | None:
    """What ties a message's fragments together: the TAG group id (a number: leading zeros name
    the same group) with the source, the first of each among the line's TAG blocks, when the line
    has a group; else the sentence's talker and id, channel and sequential message id. None when
    it is longer than KEY_CAPACITY."""
    params = [p for block in line.tag_blocks for p in block.params] if isinstance(line, Tagged) else []
    group = next((value for code, value in params if code == "g"), None)
    if group is not None:
        source = next((value for code, value in params if code == "s"), "")
        key: tuple[str, ...] = ("g", source, group.rsplit("-", 1)[-1].lstrip("0") or "0")
    else:
        # the sequential id as the fixed assemblers keep it: whether there is one, and its value
        sequence = "\0\0" if fragment.sequence is None else "\1" + chr(fragment.sequence)
        key = ("a", getattr(sentence, "talker", ""), sentence.SENTENCE, fragment.channel or "", sequence)
    return key if sum(len(part) + 1 for part in key) <= KEY_CAPACITY else None  # each part NUL-ended
