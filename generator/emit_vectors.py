"""Language-neutral test vectors: every example of the manuals, with the JSON each tool must print."""

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


def emit(spec: Spec, env: jinja2.Environment) -> dict[str, str]:
    lines = [json.dumps(v, ensure_ascii=True, separators=(",", ":")) for v in example_vectors(spec)]
    return {"vectors/examples.jsonl": "".join(line + "\n" for line in lines)}
