"""Parsing any line into the class of its sentence, and the tools' JSON in both directions."""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from typing import Any

from . import runtime
from .runtime import NmeaError
from .sentences import LAYOUTS


@dataclass(slots=True)
class Generic:
    """A well-formed sentence the spec does not describe: its address and raw fields."""

    address: str
    fields: list[str] = field(default_factory=list)
    start: str = "$"
    checksum: str | None = "upper"

    SENTENCE = None
    VARIANT = None

    def to_sentence(self) -> str:
        return runtime.assemble(self.start, self.address, self.fields, self.checksum)


def parse(line: str | bytes) -> Any:
    """Decode one sentence (a trailing CR LF is allowed) into the class of its layout, or a
    Generic for a well-formed sentence the spec does not describe. Raises NmeaError."""
    if isinstance(line, bytes):
        line = line.decode("latin-1")
    if line.endswith("\n"):
        line = line[:-2] if line.endswith("\r\n") else line[:-1]
    frame = runtime.frame(line)
    checksum = runtime.checksum_case(frame.checksum)
    address = frame.address
    layouts = LAYOUTS.get(address[2:]) if runtime.is_standard_address(frame.start, address) else None
    if layouts is None:
        return Generic(address, frame.fields, frame.start, checksum)
    first_error = None
    for layout in layouts:
        try:
            return layout.parse_fields(address[:2], frame.fields, checksum)
        except NmeaError as err:
            if first_error is None:
                first_error = err
    assert first_error is not None
    raise first_error


def to_json(sentence: Any, values: bool = False) -> str:
    """The tools' JSON line for a decoded sentence (`values`: decoded values, not texts)."""
    if isinstance(sentence, Generic):
        fields = "[" + ",".join(runtime.json_str(f) for f in sentence.fields) + "]"
        head = (f'{{"ok":true,"start":{runtime.json_str(sentence.start)},"address":{runtime.json_str(sentence.address)},'
                '"talker":null,"sentence":null,"variant":null,"fields":')
    else:
        address = sentence.talker + sentence.SENTENCE
        fields = sentence.fields_json(values)
        head = (f'{{"ok":true,"start":"$","address":{runtime.json_str(address)},"talker":{runtime.json_str(sentence.talker)},'
                f'"sentence":"{sentence.SENTENCE}","variant":{runtime.json_opt(sentence.VARIANT)},"fields":')
    text = sentence.to_sentence()
    star = text.rfind("*") if sentence.checksum is not None else -1
    checksum = runtime.json_opt(text[star + 1:] if star >= 0 else None)
    return f'{head}{fields},"checksum":{checksum}}}'


def decode_json(line: str | bytes, values: bool = False) -> str:
    """`decode`'s output for one line: the sentence as JSON, or the error as JSON."""
    try:
        return to_json(parse(line), values)
    except NmeaError as err:
        return err.to_json()


def from_json(obj: Any) -> Any:
    """Rebuild a sentence from one object of `decode`'s lossless JSON; raises NmeaError."""
    if not isinstance(obj, dict):
        raise runtime.bad_json("not a JSON object")
    checksum = runtime.checksum_case(runtime.json_opt_text(obj, "checksum"))
    sentence_id = runtime.json_opt_text(obj, "sentence")
    if sentence_id is None:
        fields = runtime.json_list(obj, "fields")
        return Generic(runtime.json_str_member(obj, "address"), [runtime.json_text(f) for f in fields],
                       runtime.json_str_member(obj, "start"), checksum)
    variant = runtime.json_opt_text(obj, "variant")
    layout = next((lay for lay in LAYOUTS.get(sentence_id, ()) if lay.VARIANT == variant), None)
    if layout is None:
        raise runtime.bad_json(f'unknown sentence "{sentence_id}"')
    fields = runtime.json_member(obj, "fields")
    if not isinstance(fields, dict):
        raise runtime.bad_json('"fields" is not an object')
    return layout.parse_fields(runtime.json_str_member(obj, "talker"), layout.fields_from_json(fields), checksum)


def encode_json(line: str) -> str:
    """`encode`'s output for one line of `decode` output: the sentence, or the error as JSON."""
    try:
        obj = json.loads(line)
    except ValueError:
        return runtime.bad_json("not JSON").to_json()
    try:
        return from_json(obj).to_sentence()
    except NmeaError as err:
        return err.to_json()
