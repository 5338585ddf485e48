"""Upgrades a spec tree written for an older schema to today's, so that `diff` and the changelog
can compare a release's spec with the working tree's (and a user's overlay written for an older
release still loads there).

Each step names the schema change it undoes, says what an old file meant in today's terms, and
leaves files already in today's form alone. The tree is rewritten in place: call it on a copy.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

import yaml

Doc = dict[str, Any]


def _manuals_maker(doc: Doc) -> bool:
    """0.1.0 named the company that makes a manual's receivers `vendor`; it is `maker` since
    "vendor" came to mean a proprietary sentence's receiver family (21026c7f)."""
    changed = False
    for entry in [*(doc.get("manuals") or []), *(doc.get("generic") or [])]:   # the generic list too
        if isinstance(entry, dict) and "vendor" in entry and "maker" not in entry:
            entry["maker"] = entry.pop("vendor")
            changed = True
    return changed


def _enum_codes(doc: Doc) -> bool:
    """Every enum says since 1a1ccd46 whether a code it does not list is kept (`open`) or refused
    (`closed`); before, every enum kept such a code, as an open one does."""
    if "enum" in doc and "codes" not in doc:
        doc["codes"] = "open"
        return True
    return False


# (the files a step reads, relative to the spec directory, and the step)
STEPS: list[tuple[str, Callable[[Doc], bool]]] = [
    ("manuals.yaml", _manuals_maker),
    ("enums/*.yaml", _enum_codes),
]


def upgrade_tree(spec: Path, *, write: bool = True) -> list[Path]:
    """The files of the spec directory `spec` that an older schema wrote, rewritten in today's
    form unless `write` is false (then only found)."""
    changed: list[Path] = []
    for pattern, step in STEPS:
        for path in sorted(spec.glob(pattern)):
            doc = yaml.safe_load(path.read_text(encoding="utf-8"))
            if isinstance(doc, dict) and step(doc):
                if write:
                    path.write_text(yaml.safe_dump(doc, sort_keys=False, allow_unicode=True), encoding="utf-8")
                changed.append(path)
    return changed
