"""Reads the spec's YAML files, keeping the line of every node, and checks them against the schema."""

from __future__ import annotations

import hashlib
import json
import pickle
import sys
from dataclasses import dataclass, field
from importlib import metadata
from pathlib import Path
from typing import Any

import jsonschema
import referencing
import yaml

from . import cache
from .errors import SpecError
from .paths import ROOT

SCHEMA_DIR = ROOT / "spec" / "schema"

Path_ = tuple[str | int, ...]


@dataclass
class Document:
    """One YAML file: its data as plain Python values, and the line of each YAML path."""

    path: Path
    data: Any
    lines: dict[Path_, int] = field(default_factory=dict)
    digest: str = ""           # of the file's text: the same text validates the same way

    def line(self, where: Path_) -> int:
        """The line of `where`, or of its nearest ancestor that has one."""
        while where not in self.lines and where:
            where = where[:-1]
        return self.lines.get(where, 1)

    def error(self, where: Path_, message: str, rule: str) -> SpecError:
        return SpecError(str(self.path), self.line(where), yaml_path(where), message, rule)


def yaml_path(where: Path_) -> str:
    out = ""
    for part in where:
        out += f"[{part}]" if isinstance(part, int) else (f".{part}" if out else part)
    return out or "(top)"


def _record_lines(node: yaml.Node, where: Path_, lines: dict[Path_, int]) -> None:
    """Remember the line of every YAML path."""
    lines[where] = node.start_mark.line + 1
    if isinstance(node, yaml.MappingNode):
        for key_node, value_node in node.value:
            _record_lines(value_node, where + (str(key_node.value),), lines)
    elif isinstance(node, yaml.SequenceNode):
        for i, item in enumerate(node.value):
            _record_lines(item, where + (i,), lines)


# libyaml's parser when PyYAML was built with it (the wheels are): the same documents, faster.
_LOADER = getattr(yaml, "CSafeLoader", yaml.SafeLoader)


# The documents parsed, by the digest of their text, pickled (a copy loads several times faster
# than YAML parses); on disk, per Python and PyYAML version.
_PARSED: dict[str, bytes] = {}
_PARSED_DIR = cache.CACHE / f"parsed-py{sys.version_info[0]}.{sys.version_info[1]}-yaml{yaml.__version__}" if cache.CACHE else None


def _parsed(digest: str) -> bytes | None:
    if digest not in _PARSED and _PARSED_DIR is not None:
        try:
            _PARSED[digest] = (_PARSED_DIR / digest).read_bytes()
        except OSError:
            return None
    return _PARSED.get(digest)


def load_document(path: Path) -> Document:
    text = path.read_text(encoding="utf-8")
    digest = hashlib.sha256(text.encode()).hexdigest()
    cached = _parsed(digest)
    if cached is not None:
        data, lines = pickle.loads(cached)
        return Document(path, data, lines, digest)
    loader = _LOADER(text)
    try:  # parsed once: the nodes give the lines, the data is built from them
        node = loader.get_single_node()
        data = loader.construct_document(node) if node is not None else None
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        raise SpecError(str(path), (mark.line + 1) if mark else 1, "(top)", f"not valid YAML: {exc}",
                        "yaml") from None
    finally:
        loader.dispose()
    lines: dict[Path_, int] = {}
    if node is not None:
        _record_lines(node, (), lines)
    _PARSED[digest] = pickle.dumps((data, lines), pickle.HIGHEST_PROTOCOL)
    if _PARSED_DIR is not None:
        cache.write_atomically(_PARSED_DIR / digest, _PARSED[digest])
    return Document(path, data, lines, digest)


_VALIDATORS: dict[str, jsonschema.Draft202012Validator] = {}
# "schema digest-of-document" of the documents found valid; on disk, one file per set of schemas
# and versions of the validating libraries, one line per document (appended by each run).
_VALID: set[str] = set()
_VALID_FILE: Path | None = None


def _validator(schema_name: str) -> jsonschema.Draft202012Validator:
    """The validator of spec/schema/`schema_name`; the schemas know each other by their $id (an
    overlay's extension refers to parts of the sentence schema)."""
    global _VALID_FILE
    if not _VALIDATORS:
        texts = {path.name: path.read_text(encoding="utf-8") for path in sorted(SCHEMA_DIR.glob("*.schema.json"))}
        schemas = {name: json.loads(text) for name, text in texts.items()}
        registry = referencing.Registry().with_resources(
            (name, referencing.Resource.from_contents(schema)) for name, schema in schemas.items())
        _VALIDATORS.update((name, jsonschema.Draft202012Validator(schema, registry=registry))
                           for name, schema in schemas.items())
        if cache.CACHE is not None:
            versions = [metadata.version(name) for name in ("jsonschema", "jsonschema-specifications", "referencing")]
            key = hashlib.sha256(json.dumps([versions, texts]).encode()).hexdigest()
            _VALID_FILE = cache.CACHE / f"valid-{key[:32]}"
            try:
                _VALID.update(_VALID_FILE.read_text(encoding="ascii").split("\n"))
            except (OSError, UnicodeDecodeError):
                pass
    return _VALIDATORS[schema_name]


def _remember_valid(entry: str) -> None:
    _VALID.add(entry)
    if _VALID_FILE is not None:
        try:  # one short line appended at once: runs side by side do not mix their lines
            _VALID_FILE.parent.mkdir(parents=True, exist_ok=True)
            with open(_VALID_FILE, "a", encoding="ascii") as out:
                out.write(entry + "\n")
        except OSError:
            pass


def schema_errors(doc: Document, schema_name: str) -> list[SpecError]:
    """Every place where `doc` breaks the JSON Schema `schema_name`."""
    validator = _validator(schema_name)
    entry = f"{schema_name} {doc.digest}"
    if doc.digest and entry in _VALID:
        return []
    errors = []
    for err in sorted(validator.iter_errors(doc.data), key=lambda e: (list(map(str, e.absolute_path)), e.message)):
        where = tuple(err.absolute_path)
        errors.append(doc.error(where, _schema_message(err), "schema"))
    if not errors and doc.digest:
        _remember_valid(entry)
    return errors


def _schema_message(err: jsonschema.ValidationError) -> str:
    """The schema's complaint; for a value that fits none of several shapes (a field or a group),
    the complaint of the shape it is closest to."""
    if err.validator == "oneOf" and err.context:
        shape = "group" if isinstance(err.instance, dict) and "group" in err.instance else None
        options = err.schema.get("oneOf", []) if isinstance(err.schema, dict) else []

        def is_group_branch(e: jsonschema.ValidationError) -> bool:
            index = e.relative_schema_path[0] if e.relative_schema_path else None
            return isinstance(index, int) and index < len(options) and "group" in str(options[index])

        branch = [e for e in err.context if (shape == "group") == is_group_branch(e)]
        best = jsonschema.exceptions.best_match(branch or err.context)
        if best is not None:
            where = "".join(f"[{p}]" if isinstance(p, int) else f".{p}" for p in best.relative_path)
            return f"{best.message}{f' (at {where[1:]})' if where else ''}"
    return err.message
