"""atheris (coverage-guided) fuzz target for the generated Python package.

Each input is tried as an NMEA line, as a line of decode's JSON, and as a byte stream cut into
chunks of sizes taken from the input itself:
- a line that parses serializes back to exactly its bytes, its JSON rebuilds the same sentence,
  and lenient parsing of it agrees; a line that does not parse raises NmeaError, nothing else;
- JSON either rebuilds a sentence that parses again, or is refused with NmeaError;
- framing a stream (binary frames too) gives the same items however it is chunked, and they
  concatenate to the stream less the line endings outside its frames.

Usage: python fuzz/python/fuzz_nmea.py [libFuzzer flags] CORPUS_DIR... (PYTHONPATH=generated/python)
"""

from __future__ import annotations

import sys

import atheris

with atheris.instrument_imports():
    import nmeaspec
    from nmeaspec import stream


def as_line(data: bytes) -> None:
    try:
        sentence = nmeaspec.parse(data)
    except nmeaspec.NmeaError:
        return
    line = data.decode("latin-1")
    if line.endswith("\n"):  # parse() takes one line ending
        line = line[:-2] if line.endswith("\r\n") else line[:-1]
    if sentence.to_sentence() != line:
        raise AssertionError(f"round trip changed {line!r} into {sentence.to_sentence()!r}")
    text = nmeaspec.to_json(sentence)
    nmeaspec.to_json(sentence, values=True)
    if nmeaspec.encode_json(text) != line:
        raise AssertionError(f"JSON round trip changed {line!r}")
    if nmeaspec.to_json(nmeaspec.parse(line, lenient=True)) != text:
        raise AssertionError(f"lenient parsing disagrees on a valid line {line!r}")


def as_json(data: bytes) -> None:
    out = nmeaspec.encode_json(data.decode("latin-1"))
    if out.startswith('{"ok":false'):
        return
    nmeaspec.parse(out)  # a rebuilt sentence must parse again (raises if it does not)


def as_stream(data: bytes) -> None:
    whole = list(stream.lines([data], binary=True))
    chunks, rest, size = [], data, 1
    while rest:
        chunks.append(rest[:size])
        rest = rest[size:]
        size = size % 7 + 1
    if list(stream.lines(chunks, binary=True)) != whole:
        raise AssertionError("framing depends on how the stream is chunked")
    if any(isinstance(item, int) for item in whole):
        return  # an overlong line's bytes are not kept
    expected, pos = bytearray(), 0
    for item in whole:
        if isinstance(item, stream.BinaryFrame):
            at = data.index(item.data, pos)
            expected += data[pos:at].replace(b"\r", b"").replace(b"\n", b"") + item.data
            pos = at + len(item.data)
    expected += data[pos:].replace(b"\r", b"").replace(b"\n", b"")
    if b"".join(item if isinstance(item, bytes) else item.data for item in whole) != expected:
        raise AssertionError("the items do not concatenate to the stream less its line endings")


def test_one_input(data: bytes) -> None:
    as_line(data)
    as_json(data)
    as_stream(data)


if __name__ == "__main__":
    atheris.Setup(sys.argv, test_one_input)
    atheris.Fuzz()
