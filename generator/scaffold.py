"""`new manual|sentence|command`: the starting YAML of a receiver's own spec files, valid as written.

A new sentence or command has one placeholder field and one example whose checksum is right, so
that `validate --spec-extra DIR` passes at once; the user then replaces the placeholders with what
the manual says, example by example.
"""

from __future__ import annotations

import re
from pathlib import Path

from .model import Spec
from .reference import rt


class ScaffoldError(ValueError):
    pass


def manual_entry(manual_id: str, maker: str, title: str) -> str:
    return f"""  - id: {manual_id}
    title: {title}
    maker: {maker}
"""


MANUALS_HEADER = """\
# The sources of this overlay's sentences and commands (the ids their `manuals:` name); laid over
# the built-in spec's manuals.yaml.
manuals:
"""


def sentence(spec: Spec, sentence_id: str, manual: str, kind: str, address: str | None) -> str:
    """A proprietary sentence (`kind` output) or command of `manual`'s receiver."""
    if not re.fullmatch(r"[A-Z][A-Z0-9_]{1,31}", sentence_id):
        raise ScaffoldError(f"{sentence_id!r} is not a sentence id: upper case letters, digits and _ (e.g. PACMEPOS)")
    address = address or sentence_id
    if not re.fullmatch(r"[A-Za-z0-9]{1,24}", address):
        raise ScaffoldError(f"give --address: {address!r} is not an address (letters and digits after $)")
    if spec.manual(manual) is None:
        raise ScaffoldError(f"unknown manual {manual!r}: add it first (`nmeaspec-gen new manual {manual} ...`)")
    existing = spec.sentence(sentence_id)
    if existing is not None:
        raise ScaffoldError(f"{sentence_id} is already defined in {existing.source}")
    body = f"{address},1"
    line = f"${body}*{rt.checksum(body):02X}"
    what = "a command the host sends" if kind == "command" else "a sentence the receiver sends"
    return f"""\
# {sentence_id}: {what} ({manual}). Replace the placeholders (name, doc, the field, the example)
# with what the manual says; `nmeaspec-gen validate --spec-extra DIR` checks the file.
sentence: {sentence_id}
address: {address}
kind: {kind}
vendor: {manual}
name: {sentence_id} {"command" if kind == "command" else "sentence"}
doc: What {sentence_id} carries, in the manual's words.
manuals: [{manual}]
fields:                            # in wire order (spec/README.md: field keys and types)
- id: value
  name: Value
  type: integer
  doc: The first field after the address.
examples:                          # the manual's example lines, verbatim, with the values they decode to
- manual: {manual}
  where: the manual's section or page
  raw: {line}
  expect: {{value: 1}}
"""


def sentence_path(overlay: Path, sentence_id: str) -> Path:
    return overlay / "proprietary" / f"{sentence_id.lower()}.yaml"
