"""Language-neutral test vectors: every example of the manuals, with the JSON each tool must print,
lines outside what the manuals allow, with what each tool prints for them by its options, and the
fixes an assembler makes of the streams of spec/fix.yaml."""

from __future__ import annotations

import json

import jinja2

from . import reference
from .model import Spec


def example_vectors(spec: Spec) -> list[dict]:
    out = []
    for sentence in spec.sentences:
        for example in sentence.examples:
            manual = spec.manual(example.manual)
            line = example.line
            record: dict = {
                "manual": manual.file if manual and manual.file else example.manual,
                "manual_id": example.manual,
                "sentence": sentence.id,
                "where": example.where,
                "raw": example.raw,
                "checksum_ok": example.checksum_ok,
                "line": line,
            }
            if example.corrected:
                record["reason"] = example.reason
            if example.unrecoverable:
                record["unrecoverable"] = example.unrecoverable
            if line is not None:
                decoded = reference.decode(spec, line)
                assert decoded.layout is not None
                record["variant"] = decoded.layout.id
                record["expect"] = json.loads(reference.expect_json(decoded.layout, example.expect or {})[0])
                record["decode"] = reference.to_json(decoded)
                record["decode_values"] = reference.to_json(decoded, values=True)
            if line != example.raw:
                # As the tools read it: the text's UTF-8 bytes, one character a byte.
                record["raw_decode"] = reference.decode_json(spec, example.raw.encode("utf-8").decode("latin-1"))
            out.append(record)
    return out


# Lines that show how parsing treats a value outside what the manual allows, each decoded with
# the tools' options below: a number outside its range is kept and flagged unless --strict; an
# unknown code of a closed enum, or a line that a variant is not there for, is refused.
TOLERANCE_LINES = (
    "$PUBX,03,02,1,-,014,-1,08,000,12,U,207,-2,28,009*5C",  # u-blox: satellites below the horizon
    "$GPRMC,225446,A,4916.45,N,12311.12,W,000.5,454.7,191194,020.3,E*6C",  # course over 359.9
    "$GPRMC,225446,X,4916.45,N,12311.12,W,000.5,054.7,191194,020.3,E*71",  # status X: closed A/V
    "$GPRMC,225446,A,4916.45,Q,12311.12,W,000.5,054.7,191194,020.3,E*77",  # hemisphere Q: not `sentinel`
)
TOLERANCE_OPTIONS = ((), ("--strict",), ("--lenient", "--strict"))


def tolerance_vectors(spec: Spec) -> list[dict]:
    return [{"line": line, "options": list(options),
             "decode": reference.decode_json(spec, line, lenient="--lenient" in options, strict="--strict" in options)}
            for line in TOLERANCE_LINES for options in TOLERANCE_OPTIONS]


def fix_vectors(spec: Spec) -> list[dict]:
    """The examples of spec/fix.yaml: lines and the facts of each fix an assembler makes of them."""
    return [{"where": e.where, "lines": e.lines, "fixes": e.expect} for e in spec.fix_examples]


def emit(spec: Spec, env: jinja2.Environment) -> dict[str, str]:
    def jsonl(records: list[dict]) -> str:
        return "".join(json.dumps(r, ensure_ascii=True, separators=(",", ":")) + "\n" for r in records)

    return {"vectors/examples.jsonl": jsonl(example_vectors(spec)),
            "vectors/tolerance.jsonl": jsonl(tolerance_vectors(spec)),
            "vectors/fixes.jsonl": jsonl(fix_vectors(spec))}
